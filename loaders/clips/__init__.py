"""Clips: time windows of a recorded log copied as raw MCAP, one pass for all windows."""

from loaders.clips.cut import MapAttachment, write_clips
from loaders.clips.errors import ClipWriteError
from loaders.clips.events import EVENT_TOPIC
from loaders.clips.model import ClipOutcome, ClipRequest
from loaders.clips.ros1_bag import write_ros1_bag

__all__ = [
    "EVENT_TOPIC",
    "ClipOutcome",
    "ClipRequest",
    "ClipWriteError",
    "MapAttachment",
    "write_clips",
    "write_ros1_bag",
]
