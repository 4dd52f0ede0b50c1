"""A drive written by ``write_drive_mcap`` reads back as the same frames and verdicts."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import pytest
from mcap.reader import make_reader

from loaders import open_drive
from loaders.records import ActorTable, EgoState, Frame
from tests.loaders.test_commonroad import basic, write
from tests.workbench.samples.drive_compare import (
    assert_same_frames,
    assert_same_verdicts,
    ego_size_of,
    verdict_records,
)
from workbench.driver import EgoSize
from workbench.drives import parse_ego_size
from workbench.errors import WorkbenchError
from workbench.samples.drive_mcap import (
    DRIVE_TOPICS,
    ego_size_option,
    frames_as_messages,
    write_drive_mcap,
)

if TYPE_CHECKING:
    from pathlib import Path


@pytest.mark.parametrize("version", ["2018b", "2020a"])
def test_commonroad_drive_reads_back_with_its_map(tmp_path: Path, version: str) -> None:
    xml = write(tmp_path, version, basic(version))
    log = tmp_path / "drive.mcap"
    source = open_drive(xml)
    assert write_drive_mcap(source, log, map_name=xml.name) == 5
    expected = list(source.frames())
    drive = open_drive(log, map=xml)
    assert drive.info.roles.ego == "/ego/odom"
    assert drive.info.roles.objects == ("/perception/objects",)
    assert drive.info.roles.plan == "/planning/trajectory"
    assert drive.lane_map is not None
    assert source.lane_map is not None
    assert len(drive.lane_map) == len(source.lane_map) == 3
    got = list(drive.frames())
    assert_same_frames(expected, got)
    # the truck, the pedestrian and the parked (unknown) vehicle keep their classes
    assert {int(c) for f in got for c in f.actors.object_class} == {0, 2, 6}
    size = ego_size_of(expected[0])
    assert_same_verdicts(verdict_records(drive, size), verdict_records(source, size))


def test_metadata_names_the_source_and_the_map(tmp_path: Path) -> None:
    xml = write(tmp_path, "2020a", basic("2020a"))
    log = tmp_path / "drive.mcap"
    write_drive_mcap(open_drive(xml), log, map_name=xml.name)
    with log.open("rb") as stream:
        reader = make_reader(stream)
        meta = {m.name: m.metadata for m in reader.iter_metadata()}
        summary = reader.get_summary()
    assert summary is not None
    topics = {c.topic: summary.schemas[c.schema_id].name for c in summary.channels.values()}
    assert topics == DRIVE_TOPICS
    assert meta["drive"]["map"] == xml.name
    assert meta["drive"]["source_ego_id"] == "10"
    assert meta["drive"]["source_format"] == "commonroad-2020a"


def test_window_limits_the_frames(tmp_path: Path) -> None:
    xml = write(tmp_path, "2020a", basic("2020a"))
    log = tmp_path / "drive.mcap"
    written = write_drive_mcap(open_drive(xml), log, window=(100_000_000, 300_000_000))
    assert written == 2
    assert [f.t_ns for f in open_drive(log, map=xml).frames()] == [100_000_000, 200_000_000]


def test_the_ego_size_option_gives_the_size_back() -> None:
    ego = EgoState(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, length_m=4.3, width_m=1.7, height_m=1.5)
    assert parse_ego_size(ego_size_option(ego)) == EgoSize(4.3, 1.7, 1.5)


def _frame(object_id: str) -> Frame:
    ego = EgoState(0.0, 0.0, 0.0, 0.0, 5.0, 0.0, 0.0)
    one = np.ones(1)
    actors = ActorTable.from_columns(
        ids=[object_id],
        object_class=[1],
        x_m=one,
        y_m=one,
        yaw_rad=one,
        vx_mps=one,
        vy_mps=one,
        length_m=one,
        width_m=one,
    )
    return Frame(3, 300, ego, actors)


@pytest.mark.parametrize("object_id", ["car7", "-1", str(2**32)])
def test_object_id_the_message_cannot_hold_is_a_one_line_error(object_id: str) -> None:
    with pytest.raises(WorkbenchError, match=rf"frame 3 \(t=300 ns\): object id '{object_id}'"):
        list(frames_as_messages([_frame(object_id)]))


def test_frame_without_plan_gets_an_empty_trajectory() -> None:
    messages = list(frames_as_messages([_frame("7")]))
    assert [topic for topic, _, _ in messages] == list(DRIVE_TOPICS)
    assert [t for _, t, _ in messages] == [300, 300, 300]
    assert messages[1][2].points == []
    assert [o.id for o in messages[0][2].objects] == [7]
