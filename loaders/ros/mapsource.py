"""Find and read the lane map of a ROS/MCAP log.

Order: ``--map FILE``; an MCAP attachment whose name ends in ``.osm``; a ``.osm`` file
beside the log with the same stem (``drive.mcap`` → ``drive.osm``); ``map.osm`` inside a
rosbag2 directory. No map is not an error (``lane_map`` is None).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from loaders.errors import MapError

if TYPE_CHECKING:
    from pathlib import Path

    from loaders.maps.model import LaneMap
    from loaders.ros.source import MessageSource

__all__ = ["find_map", "read_map"]


def read_map(source: Path | bytes, name: str) -> LaneMap:
    """Read a Lanelet2 map from a path or bytes (``name`` labels it in errors)."""
    from loaders.maps.lanelet2 import read_lanelet2  # noqa: PLC0415 - optional reader, loaded on demand

    if not isinstance(source, bytes) and source.suffix.lower() != ".osm":
        raise MapError(source, "only Lanelet2 .osm maps can accompany a ROS/MCAP log")
    return read_lanelet2(source, name=name)


def _sidecars(path: Path) -> list[Path]:
    if path.is_dir():
        return [path / "map.osm", path.with_suffix(".osm")]
    return [path.with_suffix(".osm")]


def find_map(
    path: Path, source: MessageSource, explicit: Path | None
) -> tuple[str, LaneMap] | None:
    """Return ``(description, map)`` for the log at ``path``, or None when it has none."""
    if explicit is not None:
        if not explicit.is_file():
            raise MapError(explicit, "no such map file")
        return str(explicit), read_map(explicit, str(explicit))
    for name, data in source.attachments():
        return f"attachment {name}", read_map(data, f"{path}#{name}")
    for candidate in _sidecars(path):
        if candidate.is_file():
            return str(candidate), read_map(candidate, str(candidate))
    return None
