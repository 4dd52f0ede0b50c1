"""Message logs: timestamped messages on topics (ROS 1 bags, rosbag2 directories, MCAP files).

Container sources (``rosbags_source`` for everything rosbags reads, ``mcap_source`` for MCAP
with ``ros1``/``json``/``protobuf`` channels, service-event channels or a damaged summary),
decoders per message family (``decoders``: ROS, Foxglove protobuf, our JSON), topic roles
and frame assembly on the ego clock. Not ROS-specific: an MCAP file with only Foxglove or
JSON channels is read here too.
"""

from loaders.message_logs.log_drive import LogDrive
from loaders.message_logs.registry import FAMILIES, MessageFamily

__all__ = ["FAMILIES", "LogDrive", "MessageFamily"]
