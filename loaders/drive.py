"""The ``Drive`` abstraction every reader implements."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Protocol

from loaders.timebase import ns_to_s

if TYPE_CHECKING:
    from collections.abc import Iterator
    from pathlib import Path

    from loaders.maps.model import LaneMap
    from loaders.records import Frame

__all__ = ["Drive", "DriveInfo", "TopicInfo", "TopicRoles"]


@dataclass(frozen=True, slots=True)
class TopicInfo:
    """One topic of a log."""

    topic: str
    msgtype: str
    count: int
    role: str | None = None


@dataclass(frozen=True, slots=True)
class TopicRoles:
    """Which topics feed the ego state, the actor table and the plan.

    Attributes:
        ego: The ego topic.
        objects: The object topics.
        plan: The plan topic, if any.
        ego_candidates: Every topic that could be the ego, best first (detection order).
        ego_rule: Why ``ego`` was chosen (``--ego-topic``, the profile, or the rule that
            decided among the candidates).
    """

    ego: str
    objects: tuple[str, ...] = ()
    plan: str | None = None
    ego_candidates: tuple[str, ...] = ()
    ego_rule: str = ""


@dataclass(frozen=True, slots=True)
class DriveInfo:
    """What was detected about a drive; printed by ``workbench info`` and logged as properties.

    Attributes:
        path: The drive file or bag directory.
        source_format: e.g. ``ros2-mcap``, ``ros1-mcap``, ``ros1-bag``, ``rosbag2-sqlite3``,
            ``rosbag2-mcap``,
            ``mcap-json``, ``mcap-protobuf``, ``commonroad-2020a``, ``scenario-architect``.
        start_ns: First message time.
        end_ns: Last message time.
        topics: Every topic with its type, count and detected role.
        roles: The roles in use.
        clock: Which stamp frames are built on (``log_time`` or ``header``).
        match_tolerance_ns: Objects older than this (relative to the frame) are dropped.
        frame_count: Number of frames (ego messages), exact when the index tells it.
        map_source: Where the map came from, if any.
        notes: Free-form facts worth recording (e.g. the CommonRoad ego id).
    """

    path: Path
    source_format: str
    start_ns: int
    end_ns: int
    topics: tuple[TopicInfo, ...]
    roles: TopicRoles
    clock: str = "log_time"
    match_tolerance_ns: int = 150_000_000
    frame_count: int = 0
    map_source: str | None = None
    notes: dict[str, str] = field(default_factory=dict)

    @property
    def duration_s(self) -> float:
        """Duration between first and last message."""
        return ns_to_s(self.end_ns - self.start_ns)


class Drive(Protocol):
    """A recorded drive: metadata, an optional lane map, and a stream of frames."""

    @property
    def info(self) -> DriveInfo:
        """What was detected about the drive."""
        ...

    @property
    def lane_map(self) -> LaneMap | None:
        """The drive's lane map, if it has one (attachment, sidecar, ``--map``)."""
        ...

    def frames(self, start_ns: int | None = None, end_ns: int | None = None) -> Iterator[Frame]:
        """Yield frames in time order within ``[start_ns, end_ns)``.

        Memory stays flat in the log size. A truncated or corrupted file yields every
        readable frame and then raises ``CorruptLogError``.
        """
        ...

    def close(self) -> None:
        """Release file handles."""
        ...
