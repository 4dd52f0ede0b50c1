"""Message definitions whose names cannot become Python: a typed error, not a traceback.

rosbags compiles a log's message definitions into Python classes; its grammar admits names
Python does not (a package starting with a digit). The fuzzer found it on an MCAP schema
(``tests/fuzz/corpus/mcap-ros2``); the same holds for the definitions a ROS 1 bag carries.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import pytest
from rosbags.rosbag1 import Writer as Bag1Writer
from rosbags.typesys import get_types_from_msg
from rosbags.typesys.base import TypesysError

from loaders import open_drive
from loaders.errors import LoaderError
from loaders.typestore import check_definitions, typestore
from tests.loaders import rosmsgs

if TYPE_CHECKING:
    from pathlib import Path

_POINT = "float64 x\nfloat64 y\n"


def test_well_formed_definitions_pass_unchanged() -> None:
    types = get_types_from_msg(_POINT, "geometry_msgs/msg/Point2")
    assert check_definitions(types) is types


def test_a_package_starting_with_a_digit_is_named() -> None:
    types = get_types_from_msg(_POINT, "2d_msgs/msg/Point")
    with pytest.raises(TypesysError, match=r"type name '2d_msgs' is not a Python name"):
        check_definitions(types)


def test_a_ros1_bag_with_such_a_definition_fails_in_one_line(tmp_path: Path) -> None:
    store = typestore(1)
    msgtype = "nav_msgs/msg/Odometry"
    msgdef, md5sum = store.generate_msgdef(msgtype, ros_version=1)
    assert "MSG: geometry_msgs/Point" in msgdef
    # rosbags' grammar admits the digit in a "MSG:" header only, not in a field's type
    bad = msgdef + "=" * 80 + "\nMSG: 9eometry_msgs/Extra\nfloat64 a\n"
    path = tmp_path / "bad_names.bag"
    raw = store.serialize_ros1(rosmsgs.odometry(store, 1_000_000_000), msgtype)
    with Bag1Writer(path) as writer:
        conn = writer.add_connection("/ego/odometry", msgtype, msgdef=bad, md5sum=md5sum)
        writer.write(conn, 1_000_000_000, raw)
    with pytest.raises(LoaderError) as caught:
        open_drive(path)  # rosbags registers the definitions when the bag is opened
    text = str(caught.value)
    assert "bad_names.bag" in text
    assert "not a Python name" in text
    assert "\n" not in text
