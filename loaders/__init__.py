"""Drive loaders: file formats and message types in, ``Frame`` records out; no safety logic."""

from loaders.drive import Drive, DriveInfo, TopicInfo, TopicRoles
from loaders.errors import LoaderError
from loaders.open import LOG_SUFFIXES, is_drive_path, is_rosbag2_dir, open_drive
from loaders.records import ActorTable, EgoState, Frame, ObjectClass, Plan

__all__ = [
    "LOG_SUFFIXES",
    "ActorTable",
    "Drive",
    "DriveInfo",
    "EgoState",
    "Frame",
    "LoaderError",
    "ObjectClass",
    "Plan",
    "TopicInfo",
    "TopicRoles",
    "is_drive_path",
    "is_rosbag2_dir",
    "open_drive",
]
