"""Map discovery for ROS/MCAP logs: attachment, sidecar, ``map=FILE``, none."""

from __future__ import annotations

from contextlib import closing

import pytest

from loaders import open_drive
from loaders.errors import MapError
from tests.loaders.fixtures import (
    ODOM,
    ros_entries,
    write_mcap_json,
    write_ros2_mcap,
    write_rosbag2,
)

OSM = b"""<?xml version="1.0"?>
<osm version="0.6">
  <node id="1" lat="0" lon="0"><tag k="local_x" v="0"/><tag k="local_y" v="2"/></node>
  <node id="2" lat="0" lon="0"><tag k="local_x" v="50"/><tag k="local_y" v="2"/></node>
  <node id="3" lat="0" lon="0"><tag k="local_x" v="0"/><tag k="local_y" v="-2"/></node>
  <node id="4" lat="0" lon="0"><tag k="local_x" v="50"/><tag k="local_y" v="-2"/></node>
  <way id="10"><nd ref="1"/><nd ref="2"/><tag k="type" v="line_thin"/></way>
  <way id="11"><nd ref="3"/><nd ref="4"/><tag k="type" v="line_thin"/></way>
  <relation id="100">
    <member type="way" ref="10" role="left"/><member type="way" ref="11" role="right"/>
    <tag k="type" v="lanelet"/><tag k="subtype" v="road"/>
  </relation>
</osm>
"""

CARLA = "derived_object_msgs/msg/ObjectArray"


def test_attachment(tmp_path):
    path = write_ros2_mcap(
        tmp_path / "att.mcap", ros_entries(2, ODOM, CARLA, None), attachments={"maps/town.osm": OSM}
    )
    with closing(open_drive(path)) as drive:
        assert drive.info.map_source == "attachment maps/town.osm"
        assert drive.lane_map is not None
        assert len(drive.lane_map.lanes) == 1


def test_sidecar_and_explicit_map(tmp_path):
    path = write_mcap_json(tmp_path / "drive.mcap")
    with closing(open_drive(path)) as drive:
        assert drive.lane_map is None
        assert drive.info.map_source is None
    (tmp_path / "drive.osm").write_bytes(OSM)
    with closing(open_drive(path)) as drive:
        assert drive.info.map_source == str(tmp_path / "drive.osm")
        assert drive.lane_map is not None
    explicit = tmp_path / "other.osm"
    explicit.write_bytes(OSM)
    with closing(open_drive(path, map=explicit)) as drive:
        assert drive.info.map_source == str(explicit)


def test_map_osm_inside_rosbag2_dir(tmp_path):
    bag = write_rosbag2(tmp_path / "bag", ros_entries(2, ODOM, CARLA, None), "sqlite3")
    (bag / "map.osm").write_bytes(OSM)
    with closing(open_drive(bag)) as drive:
        assert drive.lane_map is not None


def test_bad_explicit_map(tmp_path):
    path = write_mcap_json(tmp_path / "drive.mcap")
    with pytest.raises(MapError):
        open_drive(path, map=tmp_path / "missing.osm")
    broken = tmp_path / "broken.osm"
    broken.write_text("<osm")
    with pytest.raises(MapError):
        open_drive(path, map=broken)


def test_explicit_opendrive_and_commonroad_maps(tmp_path, external_dir):
    path = write_mcap_json(tmp_path / "drive.mcap")
    town = external_dir / "maps" / "Town01.xodr"
    with closing(open_drive(path, map=town)) as drive:
        assert drive.lane_map is not None
        assert drive.lane_map.format == "opendrive"
        assert len(drive.lane_map) > 100
    scenario = next(iter(sorted((external_dir / "commonroad_ngsim").glob("*.xml"))))
    with closing(open_drive(path, map=scenario)) as drive:
        assert drive.lane_map is not None
        assert drive.lane_map.format == "commonroad"
        assert len(drive.lane_map) > 0


def test_unknown_map_suffix_is_named(tmp_path):
    path = write_mcap_json(tmp_path / "drive.mcap")
    odd = tmp_path / "map.shp"
    odd.write_bytes(b"x")
    with pytest.raises(MapError, match=r"unknown map format .*\.osm, \.xodr, \.xml"):
        open_drive(path, map=odd)
