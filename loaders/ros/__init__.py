"""ROS and MCAP logs: container sources, message decoders per family, frame assembly."""

from loaders.ros.log_drive import LogDrive
from loaders.ros.registry import FAMILIES, MessageFamily

__all__ = ["FAMILIES", "LogDrive", "MessageFamily"]
