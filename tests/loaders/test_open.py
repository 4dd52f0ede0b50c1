"""What ``open_drive`` accepts by path: ``LOG_SUFFIXES`` and ``is_drive_path``."""

from __future__ import annotations

import pytest

from loaders import LOG_SUFFIXES, is_drive_path, is_rosbag2_dir, open_drive
from loaders.errors import UnsupportedFormatError


def test_suffixes_are_the_drive_formats():
    assert LOG_SUFFIXES == (".mcap", ".bag", ".db3", ".osi", ".xml", ".saa", ".scn")


@pytest.mark.parametrize("name", ["a.mcap", "b.BAG", "c.xml", "d.saa", "e.scn"])
def test_files_with_a_log_suffix_are_drives(tmp_path, name):
    path = tmp_path / name
    path.write_bytes(b"x")
    assert is_drive_path(path)


def test_other_files_and_plain_directories_are_not_drives(tmp_path):
    (tmp_path / "map.osm").write_text("<osm/>")
    (tmp_path / "notes").mkdir()
    assert not is_drive_path(tmp_path / "map.osm")
    assert not is_drive_path(tmp_path / "notes")
    assert not is_drive_path(tmp_path / "missing.mcap")
    with pytest.raises(UnsupportedFormatError, match=r"expected one of \.mcap, \.bag"):
        open_drive(tmp_path / "map.osm")


def test_a_directory_with_metadata_yaml_is_a_rosbag2_drive(tmp_path):
    bag = tmp_path / "drive_rosbag2"
    bag.mkdir()
    assert not is_rosbag2_dir(bag)
    (bag / "metadata.yaml").write_text("rosbag2_bagfile_information: {}\n")
    assert is_rosbag2_dir(bag)
    assert is_drive_path(bag)
