"""The incident event written into every clip: the fields of ``foxglove.Event``.

``foxglove.Event`` is ``start_time``, ``end_time`` (inclusive) and ``metadata`` (unique
key/value pairs). Clips of ROS logs carry it as a ROS message ``foxglove_msgs/Event`` with
those fields in the log's own encoding: rosbags 0.11 refuses an MCAP file holding any
non-ROS schema (its MCAP storage reads every schema as ROS text), so a protobuf channel
would make the whole clip unreadable to rosbags. Clips of protobuf / JSON MCAP logs carry
the protobuf ``foxglove.Event`` from ``foxglove-schemas-protobuf``.
"""

from __future__ import annotations

import functools
from typing import TYPE_CHECKING

from foxglove_schemas_protobuf.Event_pb2 import Event
from mcap_protobuf.schema import build_file_descriptor_set
from rosbags.typesys import Stores, get_types_from_msg, get_typestore

if TYPE_CHECKING:
    from rosbags.typesys.store import Typestore

__all__ = ["EVENT_TOPIC", "EventCodec", "event_codec"]

#: Topic of the clip's incident event.
EVENT_TOPIC = "/workbench/incident"

_MSGTYPE = "foxglove_msgs/msg/Event"
_EVENT_MSG = """builtin_interfaces/Time start_time
builtin_interfaces/Time end_time
foxglove_msgs/KeyValuePair[] metadata
"""
_PAIR_MSG = """string key
string value
"""


@functools.cache
def _store(ros_version: int) -> Typestore:
    store = get_typestore(Stores.ROS1_NOETIC if ros_version == 1 else Stores.ROS2_HUMBLE)
    types = get_types_from_msg(_PAIR_MSG, "foxglove_msgs/msg/KeyValuePair")
    types.update(get_types_from_msg(_EVENT_MSG, _MSGTYPE))
    store.register(types)
    return store


class EventCodec:
    """Schema and serialisation of the event for one MCAP profile."""

    def __init__(self, profile: str) -> None:
        """Choose the encoding for ``profile`` (``ros1``, ``ros2``, anything else: protobuf)."""
        self.profile = profile
        if profile in {"ros1", "ros2"}:
            version = 1 if profile == "ros1" else 2
            text, digest = _store(version).generate_msgdef(_MSGTYPE, ros_version=version)
            #: Channel metadata (ROS 1: the definition's MD5, as ROS 1 tools expect).
            self.channel_metadata = {"md5sum": digest} if version == 1 else {}
            self.schema_name = "foxglove_msgs/Event" if version == 1 else _MSGTYPE
            self.schema_encoding = f"ros{version}msg"
            self.message_encoding = "ros1" if version == 1 else "cdr"
            self.schema_data = text.encode()
        else:
            self.channel_metadata = {}
            self.schema_name = "foxglove.Event"
            self.schema_encoding = "protobuf"
            self.message_encoding = "protobuf"
            self.schema_data = build_file_descriptor_set(Event).SerializeToString()

    def encode(self, start_ns: int, end_ns: int, pairs: dict[str, str]) -> bytes:
        """Serialise one event (``start_ns``/``end_ns`` inclusive, ns)."""
        if self.profile in {"ros1", "ros2"}:
            store = _store(1 if self.profile == "ros1" else 2)
            time_t = store.types["builtin_interfaces/msg/Time"]
            pair_t = store.types["foxglove_msgs/msg/KeyValuePair"]
            msg = store.types[_MSGTYPE](
                time_t(sec=start_ns // 10**9, nanosec=start_ns % 10**9),
                time_t(sec=end_ns // 10**9, nanosec=end_ns % 10**9),
                [pair_t(key=k, value=v) for k, v in pairs.items()],
            )
            if self.profile == "ros1":
                return bytes(store.serialize_ros1(msg, _MSGTYPE))
            return bytes(store.serialize_cdr(msg, _MSGTYPE))
        event = Event()
        event.start_time.FromNanoseconds(start_ns)
        event.end_time.FromNanoseconds(end_ns)
        for key, value in pairs.items():
            item = event.metadata.add()
            item.key = key
            item.value = value
        return bytes(event.SerializeToString())


@functools.cache
def event_codec(profile: str) -> EventCodec:
    """The (cached) :class:`EventCodec` of ``profile``."""
    return EventCodec(profile)
