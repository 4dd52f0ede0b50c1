"""Find and read the lane map of a ROS/MCAP log.

Order: ``--map FILE`` (Lanelet2 ``.osm``, OpenDRIVE ``.xodr`` or CommonRoad ``.xml``); an
MCAP attachment whose name ends in ``.osm``; a ``.osm`` file beside the log with the same
stem (``drive.mcap`` → ``drive.osm``); ``map.osm`` inside a rosbag2 directory. No map is
not an error (``lane_map`` is None).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from loaders.errors import MapError

if TYPE_CHECKING:
    from pathlib import Path

    from loaders.maps.model import LaneMap
    from loaders.message_logs.source import MessageSource

__all__ = ["find_map", "read_map", "sidecar_candidates", "sidecar_map"]


def read_map(source: Path | bytes, name: str) -> LaneMap:
    """Read a map from a path or bytes (``name`` labels it in errors).

    Bytes (MCAP attachments) are Lanelet2. A ``--map`` path may be Lanelet2 ``.osm``,
    OpenDRIVE ``.xodr`` or the lanelet network of a CommonRoad ``.xml``.
    """
    # Readers load on demand: most logs need one of them at most.
    from loaders.maps.commonroad import read_commonroad_map  # noqa: PLC0415
    from loaders.maps.lanelet2 import read_lanelet2  # noqa: PLC0415
    from loaders.maps.opendrive import read_opendrive  # noqa: PLC0415

    if isinstance(source, bytes):
        return read_lanelet2(source, name=name)
    readers = {".osm": read_lanelet2, ".xodr": read_opendrive, ".xml": read_commonroad_map}
    reader = readers.get(source.suffix.lower())
    if reader is None:
        known = ", ".join(readers)
        raise MapError(source, f"unknown map format (known: {known})", value=source.suffix)
    return reader(source, name=name)


def sidecar_candidates(path: Path) -> list[Path]:
    """Where a sidecar map of the log may lie, in the order they are tried (existing or not)."""
    if path.is_dir():
        return [path / "map.osm", path.with_suffix(".osm")]
    return [path.with_suffix(".osm")]


def sidecar_map(path: Path) -> Path | None:
    """The map file lying beside the log (``LOG.osm``; in a bag directory ``map.osm``), if any."""
    return next((c for c in sidecar_candidates(path) if c.is_file()), None)


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
    candidate = sidecar_map(path)
    if candidate is not None:
        return str(candidate), read_map(candidate, str(candidate))
    return None
