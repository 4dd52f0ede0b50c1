"""Every committed sample opens with its reader and carries the expected topics and counts."""

from __future__ import annotations

import json
from typing import Any

import jsonschema
import pytest
from mcap.reader import make_reader
from mcap_protobuf.decoder import DecoderFactory
from rosbags.highlevel import AnyReader

from tests.workbench.samples.conftest import SAMPLE_DIR
from workbench.samples.foxglove_writer import FOXGLOVE_TOPICS
from workbench.samples.generate import FOXGLOVE_SCENARIO, SCENARIOS
from workbench.samples.ros_writers import topic_types

VARIANTS = [("mcap", 2), ("bag", 1), ("rosbag2", 2)]


def _path(name: str, variant: str):
    return SAMPLE_DIR / (f"{name}_rosbag2" if variant == "rosbag2" else f"{name}.{variant}")


def _expected_counts(n_samples: int, types: dict[str, str]) -> dict[str, int]:
    per_10hz = (n_samples + 1) // 2
    topics = list(types)
    return {t: n_samples if i == 0 or t == "/tf" else per_10hz for i, t in enumerate(topics)}


@pytest.mark.parametrize("name", list(SCENARIOS))
@pytest.mark.parametrize(("variant", "ros_version"), VARIANTS)
def test_ros_files_open_with_anyreader(name, variant, ros_version):
    sc = SCENARIOS[name]()
    types = topic_types(sc, ros_version)
    with AnyReader([_path(name, variant)]) as reader:
        found = {c.topic: c.msgtype for c in reader.connections}
        counts = {c.topic: c.msgcount for c in reader.connections}
        assert found == types
        assert counts == _expected_counts(len(sc.t_s), types)
        seen: set[str] = set()
        for conn, t_ns, raw in reader.messages():
            if conn.topic in seen:
                continue
            seen.add(conn.topic)
            msg: Any = reader.deserialize(raw, conn.msgtype)
            stamp = msg.transforms[0].header.stamp if conn.topic == "/tf" else msg.header.stamp
            assert stamp.sec * 10**9 + stamp.nanosec == t_ns
        assert seen == set(types)


@pytest.mark.parametrize("name", list(SCENARIOS))
def test_mcap_has_map_attachment_and_drive_metadata(name):
    osm = (SAMPLE_DIR / f"{name}.osm").read_bytes()
    with (SAMPLE_DIR / f"{name}.mcap").open("rb") as stream:
        reader = make_reader(stream)
        attachments = list(reader.iter_attachments())
        metadata = {m.name: m.metadata for m in reader.iter_metadata()}
    assert [(a.name, a.media_type) for a in attachments] == [(f"{name}.osm", "application/xml")]
    assert attachments[0].data == osm
    assert metadata["drive"]["scenario"] == name
    assert metadata["drive"]["map"] == f"{name}.osm"
    assert (SAMPLE_DIR / f"{name}_rosbag2" / "map.osm").read_bytes() == osm


def test_foxglove_mcap_decodes():
    name = FOXGLOVE_SCENARIO
    sc = SCENARIOS[name]()
    counts: dict[str, int] = dict.fromkeys(FOXGLOVE_TOPICS, 0)
    with (SAMPLE_DIR / f"{name}_foxglove.mcap").open("rb") as stream:
        reader = make_reader(stream, decoder_factories=[DecoderFactory()])
        summary = reader.get_summary()
        assert summary is not None
        schemas = {ch.topic: summary.schemas[ch.schema_id].name for ch in summary.channels.values()}
        assert schemas == FOXGLOVE_TOPICS
        plan_schema = json.loads(
            next(s for s in summary.schemas.values() if s.encoding == "jsonschema").data
        )
        for _schema, channel, message in reader.iter_messages():
            counts[channel.topic] += 1
            if channel.message_encoding == "json":
                plan = json.loads(message.data)
                jsonschema.validate(plan, plan_schema)
                assert plan["t_ns"] == message.log_time
                assert len({len(plan[k]) for k in plan if k != "t_ns"}) == 1
        stream.seek(0)
        reader = make_reader(stream, decoder_factories=[DecoderFactory()])
        update = next(m for _, _, _, m in reader.iter_decoded_messages(topics=["/scene/objects"]))
        keys = {kv.key for kv in update.entities[0].metadata}
        assert keys == {"class", "vx_mps", "vy_mps"}
        assert len(update.entities[0].cubes) == 1
    assert counts == {
        "/ego/odometry": len(sc.t_s),
        "/scene/objects": (len(sc.t_s) + 1) // 2,
        "/planning/plan": (len(sc.t_s) + 1) // 2,
    }
