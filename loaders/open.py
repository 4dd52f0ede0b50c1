"""``open_drive``: one entry point choosing a reader by suffix and content.

| input                                   | reader                                   |
|-----------------------------------------|------------------------------------------|
| ``.bag``                                | rosbags ``AnyReader`` (ROS 1)            |
| rosbag2 directory (sqlite3 or mcap)     | rosbags ``AnyReader``                    |
| ``.db3`` (rosbag2 storage, no metadata) | rosbags ``AnyReader``                    |
| ``.osi`` (ASAM OSI trace, gt / sv)      | ``betterosi``                            |
| ``.mcap`` with ``cdr`` channels         | ``AnyReader`` (``mcap`` if summary damaged |
|                                         | or service-event channels present)       |
| ``.mcap`` with ``ros1``/``json``/``protobuf`` | ``mcap`` reader (OSI: ``betterosi``) |
| ``.xml`` (CommonRoad)                   | ``loaders.commonroad``                   |
| ``.saa`` / ``.scn`` (ScenarioArchitect) | ``loaders.scenario_architect``           |
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

from loaders.errors import (
    EmptyLogError,
    LoaderError,
    LogNotFoundError,
    UnsupportedFormatError,
)
from loaders.message_logs.assemble import AssemblyOptions
from loaders.message_logs.ego_streams import ego_settings
from loaders.message_logs.log_drive import LogDrive
from loaders.message_logs.mapsource import find_map, read_map
from loaders.message_logs.mcap_source import McapSource
from loaders.message_logs.osi_source import OsiTraceSource
from loaders.message_logs.roles import detect_roles
from loaders.message_logs.rosbags_source import RosbagsSource
from loaders.profile import DEFAULT_TOLERANCE_NS, Profile, load_profile

if TYPE_CHECKING:
    from loaders.drive import Drive
    from loaders.message_logs.source import MessageSource

__all__ = ["LOG_SUFFIXES", "SCENARIO_SUFFIXES", "is_drive_path", "is_rosbag2_dir", "open_drive"]

#: File suffixes ``open_drive`` accepts (lower case; besides rosbag2 directories).
LOG_SUFFIXES: tuple[str, ...] = (".mcap", ".bag", ".db3", ".osi", ".xml", ".saa", ".scn")
#: Suffixes of the drives that are not message logs (CommonRoad, ScenarioArchitect): no
#: sidecar map.
SCENARIO_SUFFIXES = frozenset({".xml", ".saa", ".scn"})


def is_rosbag2_dir(path: Path) -> bool:
    """Whether ``path`` is a rosbag2 bag: a directory holding ``metadata.yaml``."""
    return path.is_dir() and (path / "metadata.yaml").is_file()


def is_drive_path(path: Path) -> bool:
    """Whether ``path`` is a drive ``open_drive`` takes, judged by its kind only.

    A drive is a file with one of :data:`LOG_SUFFIXES` (any case) or a rosbag2 directory;
    the content is not checked.
    """
    return (path.is_file() and path.suffix.lower() in LOG_SUFFIXES) or is_rosbag2_dir(path)


def _rosbag2_storage(path: Path) -> str:
    if any(path.glob("*.db3")):
        return "rosbag2-sqlite3"
    if any(path.glob("*.mcap")):
        return "rosbag2-mcap"
    raise UnsupportedFormatError(path, "directory is not a rosbag2 bag (no .db3 or .mcap inside)")


def _open_source(path: Path) -> MessageSource:
    if path.is_dir():
        if not is_rosbag2_dir(path):
            raise UnsupportedFormatError(path, "directory without rosbag2 metadata.yaml")
        return RosbagsSource(path, _rosbag2_storage(path))
    if path.stat().st_size == 0:
        raise EmptyLogError(path, "file has 0 bytes")
    suffix = path.suffix.lower()
    if suffix == ".bag":
        return RosbagsSource(path, "ros1-bag")
    if suffix == ".db3":
        return RosbagsSource(path, "rosbag2-sqlite3")  # a bare storage file: topics table
    if suffix == ".osi":
        return OsiTraceSource(path)  # ASAM OSI trace: GroundTruth / SensorView
    source = McapSource(path)
    if source.source_format == "ros2-mcap" and source.indexed and not source.ignored:
        source.close()
        return RosbagsSource(path, "ros2-mcap")
    return source


def _profile(profile: str | Path | Profile | None) -> Profile | None:
    if profile is None or isinstance(profile, Profile):
        return profile
    return load_profile(profile)


def _open_other(
    path: Path, suffix: str, map_path: Path | None, ego_id: str | None, plan: Any
) -> Drive:
    if suffix == ".xml":
        from loaders.commonroad import open_commonroad  # noqa: PLC0415 - optional reader, loaded on demand

        lane_map = None if map_path is None else read_map(map_path, str(map_path))
        return open_commonroad(path, ego_id=ego_id, lane_map=lane_map)
    from loaders.scenario_architect import open_scenario_architect  # noqa: PLC0415 - optional reader

    return (
        open_scenario_architect(path) if plan is None else open_scenario_architect(path, plan=plan)
    )


def open_drive(
    path: str | Path,
    *,
    map: str | Path | None = None,  # noqa: A002 - mirrors the CLI option --map
    profile: str | Path | Profile | None = None,
    ego_id: str | None = None,
    window: tuple[int | None, int | None] | None = None,
    plan: str | None = None,
    ego_topic: str | None = None,
) -> Drive:
    """Open a recorded drive.

    Args:
        path: ``.mcap``, ``.bag``, rosbag2 directory, ``.db3``, ASAM OSI ``.osi``,
            CommonRoad ``.xml`` or ScenarioArchitect ``.saa``/``.scn``.
        map: Lane map file (Lanelet2 ``.osm`` for ROS/MCAP logs); default: attachment or
            sidecar file.
        profile: TOML topic profile (path or parsed ``Profile``).
        ego_id: CommonRoad obstacle promoted to ego; for ROS/MCAP logs, an object id
            removed from the actor tables (the ego's own entry in a global object list).
        window: ``(start_ns, end_ns)`` bounds of the frames ``frames()`` yields.
        plan: ScenarioArchitect trajectory used as plan (``emergency``/``performance``).
        ego_topic: The ego topic of a ROS/MCAP log (``--ego-topic``), over the profile's and
            the detected one.

    Returns:
        The drive; close it when done.

    Raises:
        LoaderError: A subclass naming the file and what is wrong with it.
    """
    path = Path(path)
    map_path = None if map is None else Path(map)
    if not path.exists():
        raise LogNotFoundError(path)
    suffix = path.suffix.lower()
    if path.is_file() and suffix not in LOG_SUFFIXES:
        raise UnsupportedFormatError(
            path, f"suffix {suffix or '(none)'}; expected one of {', '.join(LOG_SUFFIXES)}"
        )
    if suffix in SCENARIO_SUFFIXES:
        return _open_other(path, suffix, map_path, ego_id, plan)
    prof = _profile(profile)
    source = _open_source(path)
    try:
        roles = detect_roles(path, source.topics, prof, ego_topic)
        lane_map = find_map(path, source, map_path)
        ego = ego_settings(source, roles, prof, None if lane_map is None else lane_map[1])
    except LoaderError:
        source.close()
        raise
    start, end = window or (None, None)
    options = AssemblyOptions(
        clock=prof.clock if prof else "log_time",
        tolerance_ns=prof.match_tolerance_ns if prof else DEFAULT_TOLERANCE_NS,
        invalid_ego=prof.invalid_ego if prof else "raise",
        exclude_id=None if ego_id is None else str(ego_id),
        start_ns=start,
        end_ns=end,
    )
    return LogDrive(source, roles, options, lane_map, ego)
